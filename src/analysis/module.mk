# Layer: analysis. Modules and the objects of the modules each one uses.
MODULES += analysis analysis_events assembly body_elements condensed_contact condensed_equilibrium dof_numbering equilibrium \
           equilibrium_common increment_results load_state
$(OBJDIR)/analysis.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/assembly.o $(OBJDIR)/condensed_contact.o $(OBJDIR)/contact.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/equilibrium.o $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/load_state.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/analysis_events.o: $(OBJDIR)/increment_results.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/assembly.o: $(OBJDIR)/body_elements.o $(OBJDIR)/contact.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/element_library.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/body_elements.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/model.o
$(OBJDIR)/condensed_contact.o: $(OBJDIR)/assembly.o $(OBJDIR)/contact.o $(OBJDIR)/dense_cholesky.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/element_interface.o $(OBJDIR)/element_library.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/model.o $(OBJDIR)/solver_codes.o
$(OBJDIR)/dof_numbering.o: $(OBJDIR)/contact.o $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/model.o $(OBJDIR)/ordering.o
$(OBJDIR)/condensed_equilibrium.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/assembly.o $(OBJDIR)/condensed_contact.o $(OBJDIR)/contact.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/equilibrium_common.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/model.o
$(OBJDIR)/equilibrium.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/assembly.o $(OBJDIR)/condensed_equilibrium.o $(OBJDIR)/contact.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/equilibrium_common.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/messages.o $(OBJDIR)/model.o
$(OBJDIR)/equilibrium_common.o: $(OBJDIR)/analysis_events.o $(OBJDIR)/assembly.o $(OBJDIR)/condensed_contact.o $(OBJDIR)/contact.o $(OBJDIR)/dof_numbering.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/increment_results.o: $(OBJDIR)/assembly.o $(OBJDIR)/contact.o $(OBJDIR)/contact_results.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
$(OBJDIR)/load_state.o: $(OBJDIR)/assembly.o $(OBJDIR)/distributed_loads.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/strings.o
